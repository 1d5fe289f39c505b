Comment: roadbrdf regression input, hand-written
Version: 2.2
Channels: 1e30
Data:
Wvl	Reflect. %
400	50
