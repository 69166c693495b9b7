set key noenhanced  # exp_plot: titles are plain names
set datafile columnheaders  # exp_plot: each CSV block starts with a header line
set datafile separator comma
set logscale x
set grid
set xlabel 'LUT size N'
set ylabel 'ns per pixel (median)'
set key top left
set xtics (2,4,8,16,32,64)
plot 'size_curves.csv' index 12 using 3:8 with linespoints title 'trilinear', '' index 14 using 3:8 with linespoints title 'tetrahedral'
