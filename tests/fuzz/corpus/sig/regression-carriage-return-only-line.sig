/*** Spectra Vista SIG Data ***/
units= Counts, Counts
data=
400 10 5 50

410 10 5 50
