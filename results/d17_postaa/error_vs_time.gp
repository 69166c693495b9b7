set datafile separator comma
set xlabel 'ns per pixel (median)'
set ylabel 'RMS error on edge pixels'
set grid
set key off
set logscale x
set offsets graph 0.1, graph 0.3, graph 0.1, graph 0.1
plot 'error_vs_time.csv' using 2:3 with points pt 7 ps 1.5, '' using 2:3:1 with labels left rotate by 20 offset 1,0.5
