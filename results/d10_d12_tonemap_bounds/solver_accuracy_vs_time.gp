set datafile separator comma
set logscale xy
set xlabel 'ns per inverse (median)'
set ylabel 'max relative error of c'
set grid
set key outside right
set format y '10^{%L}'
plot 'solver_curves.csv' index 0 using 5:4 with linespoints title 'filmic-hbd bisection', '' index 1 using 5:4 with linespoints title 'filmic-hbd Newton', '' index 2 using 5:4 with linespoints title 'aces-fit bisection', '' index 3 using 5:4 with linespoints title 'aces-fit Newton', '' index 4 using 5:4 with linespoints title 'aces-rrt-odt bisection', '' index 5 using 5:4 with linespoints title 'aces-rrt-odt Newton'
