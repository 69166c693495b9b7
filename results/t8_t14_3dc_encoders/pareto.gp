set logscale x
set xlabel 'encode time per 4x4 block (core-ns)'
set ylabel 'RMS angular error (deg), 16-bit interpolation'
set grid
set key off
plot 'pareto.dat' using 2:3 with points pt 7 ps 1.2, '' using 2:3:1 with labels offset 0,1 font ',8'

