set key noenhanced  # exp_plot: titles are plain names
set datafile separator comma
set xlabel 'alpha'
set ylabel 'mean angular error (deg)'
set logscale y
set grid
set key outside right
plot for [c=2:4] 'blending_plot.csv' skip 1 using 1:c with linespoints lc c title 'best fit, '.word('5 30 90', c-1).' deg', for [c=5:7] '' skip 1 using 1:c with linespoints dt 2 lc (c-3) title 'normalized, '.word('5 30 90', c-4).' deg'
