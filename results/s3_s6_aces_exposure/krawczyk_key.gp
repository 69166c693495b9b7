set key noenhanced  # exp_plot: titles are plain names
set datafile columnheaders  # exp_plot: each CSV block starts with a header line
set datafile separator comma
set grid
set xlabel 'EV100'
set ylabel 'key value'
plot 'krawczyk_curve.csv' using 1:2 with lines lw 2 title '1.03 - 2/(log10(L+1)+2)'
