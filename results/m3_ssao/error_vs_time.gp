set key noenhanced  # exp_plot: titles are plain names
set datafile columnheaders  # exp_plot: each CSV block starts with a header line
set datafile separator comma
set logscale xy
set xlabel 'ns per full-resolution pixel (median)'
set ylabel 'RMS error of VO'
set grid
set key top right
plot 'samples_curves.csv' using 3:2:1 with linespoints lw 2 title 'full resolution', '' using 3:2:1 with labels offset 0,1 notitle, '' using 5:4 with linespoints title 'half resolution', '' using 5:4:1 with labels offset 0,-1 notitle
