set key noenhanced  # exp_plot: titles are plain names
set datafile separator comma
set logscale xy
set xlabel 'quadrature samples per axis'
set ylabel 'max abs error vs the finest grid'
set grid
plot 'convergence_points.csv' every ::1 using 1:2 with linespoints pt 7 title 'scale/bias'

