set key noenhanced  # exp_plot: titles are plain names
set datafile columnheaders  # exp_plot: each CSV block starts with a header line
set datafile separator comma
set key autotitle columnhead top left
set grid
set xlabel 'time (s)'
set ylabel 'EV100'
plot for [i=2:5] 'exposure_frames.csv' using 1:i with lines lw 2, '' using 1:6 with lines lw 4
