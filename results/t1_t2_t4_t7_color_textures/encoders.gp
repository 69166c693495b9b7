set key noenhanced  # exp_plot: titles are plain names
set datafile separator comma
set grid
set logscale x
set key top right
set xlabel 'ns per texel (one thread)'
set ylabel 'RMS error (8-bit units)'
plot 'encoder_points.csv' skip 1 using ($4==0?$3:1/0):2 with points pt 7 ps 1.2 title 'sol', '' skip 1 using ($4==1?$3:1/0):2 with points pt 5 ps 1.2 title 'libsquish'
