set key noenhanced  # exp_plot: titles are plain names
set datafile columnheaders  # exp_plot: each CSV block starts with a header line
set datafile separator comma
set logscale xy
set grid
set xlabel 'LUT size N'
set ylabel 'max CIEDE2000 over the 8-bit cube'
set key outside right
set xtics (2,4,8,16,32,64)
plot for [l=0:4] 'size_curves.csv' index 3*l+1 using 3:6 with linespoints title sprintf('look %d, tri 8-bit', l), for [l=0:4] '' index 3*l+2 using 3:6 with linespoints dt 2 title sprintf('look %d, tetra', l), 1 with lines lc rgb 'black' dt 3 title 'dE00 = 1'
