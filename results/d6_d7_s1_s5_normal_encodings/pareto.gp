set datafile separator comma
set logscale xy
set xlabel 'ns per normal (encode + decode)'
set ylabel 'RMS angular error (deg)'
set grid
set key off
set offsets graph 0.05, graph 0.3, 0, 0
plot 'pareto.csv' skip 1 using 2:3 with points pt 7 ps 1.2, '' skip 1 using 2:3:1 with labels offset char 1,0.5 left font ',7'
