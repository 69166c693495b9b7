set key noenhanced  # exp_plot: titles are plain names
set datafile columnheaders  # exp_plot: each CSV block starts with a header line
set datafile separator comma
set xlabel 'frame (panning camera)'
set ylabel 'RMS error vs supersampled frame'
set grid
set key top right
plot 'error_per_frame.csv' using 1:2 with lines lw 2 title 'aliased', '' using 1:3 with lines title 'post-process AA', '' using 1:4 with lines lw 2 title 'TAA (jitter + 3x3 depth test)', '' using 1:5 with lines dt 4 title 'TAA, 1-pixel depth test', '' using 1:6 with lines dt 2 title 'TAA without depth test', '' using 1:7 with lines dt 3 title 'TAA without jitter'
