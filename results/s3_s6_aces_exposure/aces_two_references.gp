set key noenhanced  # exp_plot: titles are plain names
set datafile columnheaders  # exp_plot: each CSV block starts with a header line
set datafile separator comma
set key autotitle columnhead bottom right
set grid
set xlabel 'x (scene value)'
set ylabel 'linear display value'
plot 'hill_curves.csv' using 1:2 with lines lw 2 title 'Narkowicz fit(x)', '' using 1:3 with lines lw 2 title 'Hill ACESFitted(2x)', '' using 1:4 with lines dt 2 title 'ACES 1.0 ref(2x)'
