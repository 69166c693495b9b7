set key noenhanced  # exp_plot: titles are plain names
set datafile separator comma
set logscale x 2
set logscale y
set xlabel 'table size (texels per side)'
set ylabel 'RMS angular error (deg)'
set grid
set key top right
plot 'table_sweep_plot.csv' skip 1 using 1:2 with linespoints lw 3 title '8-bit, nearest', '' skip 1 using 1:3 with linespoints title '16-bit, nearest', '' skip 1 using 1:4 with linespoints dt 3 title 'float, nearest', '' skip 1 using 1:5 with linespoints title '16-bit, bilinear', 0.036773 with lines dt 2 title 'exact search'
