set key noenhanced  # exp_plot: titles are plain names
set datafile separator comma
set logscale xy
set key outside right
set grid
set xlabel 'LUT texels per side (ns per lookup: see the table)'
set ylabel 'abs error of F0*scale+bias, F0=0.04'
set xrange [6:160]
plot 'error_vs_time.csv' every ::1 using 1:2 with linespoints pt 7 title 'LUT, max', '' every ::1 using 1:3 with linespoints pt 6 title 'LUT, mean', 0.115646 with lines dt 2 lc rgb 'red' title 'polynomial, max', 0.00901622 with lines dt 3 lc rgb 'red' title 'polynomial, mean', 0.0813193 with lines dt 2 lc rgb 'blue' title 'Lazarov refit, max', 0.0104551 with lines dt 3 lc rgb 'blue' title 'Lazarov refit, mean'

