set key noenhanced  # exp_plot: titles are plain names
set datafile columnheaders  # exp_plot: each CSV block starts with a header line
set datafile separator comma
set logscale xy
set format x '10^{%L}'
set format y '10^{%L}'
set xlabel 'x = c / l'
set ylabel 'tone-mapped linear output'
set key top left
set grid
set yrange [1e-5:1.2]
plot for [i=2:7] 'curves.csv' using 1:i with lines lw 2 title columnheader(i), 0.00196078431 with lines dt 2 lc rgb 'black' title 'LDR threshold 1/510'
