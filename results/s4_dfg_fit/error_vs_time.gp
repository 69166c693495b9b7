set datafile separator comma
set logscale xy
set key top right
set xlabel 'ns per evaluation (CPU)'
set ylabel 'max abs error, F0=0.04'
plot 'error_vs_time.csv' every ::1 using 4:2:1 with labels offset char 0,1 notitle, '' every ::1 using 4:2 with points pt 7 title 'max error', '' every ::1 using 4:3 with points pt 6 title 'mean error'

