set key noenhanced  # exp_plot: titles are plain names
set datafile columnheaders  # exp_plot: each CSV block starts with a header line
set datafile separator comma
set grid
set xlabel 'input scale s in ref(s x)'
set ylabel 'max |fit(x) - ref(s x)|, x in [0,16]'
set logscale y
plot 'scale_sweep_curve.csv' using 1:2 with lines lw 2 notitle
