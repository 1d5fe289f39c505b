Version: 2.3 [1.0.5136]
Channels: 1e30
Data:
Wvl	Reflect. %
400	50
