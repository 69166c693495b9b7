set key noenhanced  # exp_plot: titles are plain names
set datafile columnheaders  # exp_plot: each CSV block starts with a header line
set datafile separator comma
set xlabel 'frame (panning camera)'
set ylabel 'RMS error where the moving box recently was'
set grid
set key top left
plot 'error_per_frame.csv' using 1:8 with linespoints title 'TAA, 3x3 depth test', '' using 1:9 with linespoints title 'TAA, 1-pixel depth test', '' using 1:10 with linespoints title 'TAA without depth test (ghosting)'
