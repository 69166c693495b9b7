set key noenhanced  # exp_plot: titles are plain names
set datafile columnheaders  # exp_plot: each CSV block starts with a header line
set datafile separator comma
set xlabel 'test cost (ns per box, median)'
set ylabel 'hidden boxes culled (%)'
set key bottom right
set grid
plot 'refine_curves.csv' index 0 using 6:3 with linespoints lw 2 title 'max downscale (conservative)', '' index 1 using 6:3 with linespoints title 'min downscale', '' index 2 using 6:3 with linespoints title 'mean downscale'
