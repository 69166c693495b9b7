set key noenhanced  # exp_plot: titles are plain names
set logscale x
set offsets graph 0, graph 0.2, graph 0.12, graph 0.02
set xlabel 'encode time per 4x4 block (core-ns)'
set ylabel 'RMS angular error (deg), 16-bit interpolation'
set grid
set key off
plot 'pareto.dat' using 2:3 with points pt 7 ps 1.2, '' using 2:3:1 with labels rotate by 35 left offset 0.6,0.6 font ',8'

