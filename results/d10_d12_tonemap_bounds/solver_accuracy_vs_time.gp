set key noenhanced  # exp_plot: titles are plain names
set datafile columnheaders  # exp_plot: each CSV block starts with a header line
set datafile separator comma
set logscale xy
set xlabel 'ns per inverse (median)'
set ylabel 'max relative error of c'
set grid
set key outside right
set format y '10^{%L}'
set yrange [1e-17:1e-1]
plot 'solver_curves.csv' index 0 using 5:4 with linespoints title 'filmic-hbd bisection', '' index 1 using 5:4 with linespoints title 'filmic-hbd Newton', '' index 2 using 5:4 with linespoints title 'aces-fit bisection', '' index 3 using 5:4 with linespoints title 'aces-fit Newton', '' index 4 using 5:4 with linespoints title 'aces-rrt-odt bisection', '' index 5 using 5:4 with linespoints title 'aces-rrt-odt Newton', 'solver_closed_form.csv' using 2:(1e-16) with points pt 7 ps 1.5 title 'closed forms (exact; drawn at 1e-16)'
