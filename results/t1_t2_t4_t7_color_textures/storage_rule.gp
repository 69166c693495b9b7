set key noenhanced  # exp_plot: titles are plain names
set datafile separator comma
set grid
set key outside below
set xlabel 'share of values above the median'
set ylabel 'log2(RMS gamma / RMS linear)'
set arrow from 0.75,graph 0 to 0.75,graph 1 nohead dt 2 lc rgb 'gray'
set label '75%' at 0.76,graph 0.05 tc rgb 'gray'
set xzeroaxis lw 2
plot 'storage_points.csv' skip 1 using 1:3 with points pt 7 ps 0.6 title 'linear light, median 60/255', '' skip 1 using 2:3 with points pt 6 ps 0.6 title 'linear light, median 116/255', '' skip 1 using 1:4 with points pt 5 ps 0.6 title 'display after exposure, median 60/255'
