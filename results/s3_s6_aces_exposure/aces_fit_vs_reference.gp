set key noenhanced  # exp_plot: titles are plain names
set datafile columnheaders  # exp_plot: each CSV block starts with a header line
set datafile separator comma
set key autotitle columnhead bottom right
set grid
set xlabel 'x (scene value)'
set ylabel 'linear display value'
set y2label 'fit - ref(2x)'
set y2tics
set ytics nomirror
plot 'aces_curves.csv' using 1:2 with lines lw 2 title 'ACES fit', '' using 1:3 with lines lw 2 title 'RRT+ODT ref(2x)', '' using 1:4 with lines dt 2 title 'ref(x/0.6)', '' using 1:5 axes x1y2 with lines lc rgb 'red' title 'fit - ref(2x) (right axis)'
