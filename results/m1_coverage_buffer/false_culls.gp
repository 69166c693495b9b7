set key noenhanced  # exp_plot: titles are plain names
set datafile columnheaders  # exp_plot: each CSV block starts with a header line
set datafile separator comma
set style data histograms
set style fill solid 0.6
set xlabel 'refinement levels below the start level'
set ylabel 'visible boxes culled'
set grid ytics
set key top left
plot 'refine_curves.csv' index 0 using 4:xtic(2) title 'max', '' index 1 using 4 title 'min', '' index 2 using 4 title 'mean'
