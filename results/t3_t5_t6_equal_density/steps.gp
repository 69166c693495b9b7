set key noenhanced  # exp_plot: titles are plain names
set datafile columnheaders  # exp_plot: each CSV block starts with a header line
set datafile separator comma
set grid
set logscale y 2
set key top left
set xlabel 'linear value x'
set ylabel '8-bit step / linear storage step (1/255)'
set xrange [0:1]
set yrange [0.05:4]
set arrow from 5.0/11,0.05 to 5.0/11,4 nohead dt 2 lc rgb 'gray'
set label 'talk 5/11' at 5.0/11+0.01,0.08 tc rgb 'gray'
plot 'steps.csv' using 1:2 with lines lw 2 title 'linear', '' using 1:3 with lines lw 2 title 'power 2.2', '' using 1:4 with lines title 'sRGB', '' using 1:5 with steps lw 2 title 'Xbox 360 PWL'
