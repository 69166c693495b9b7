set key noenhanced  # exp_plot: titles are plain names
set datafile columnheaders  # exp_plot: each CSV block starts with a header line
set datafile separator comma
set grid
set logscale y
set format y '10^{%L}'
set yrange [1e-9:1e-2]
set xlabel 'linear depth (around x = 100/255)'
set ylabel '|decoded - depth|'
set key top left
plot 'edge_errors.csv' using 1:($2+1e-12) with lines title 'UNORM16', '' using 1:($3+1e-12) with lines lw 2 title 'x + y/255 (x = floor)', '' using 1:($4+1e-12) with lines title 'x rounded by the UNORM write'
