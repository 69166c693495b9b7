set key noenhanced  # exp_plot: titles are plain names
set datafile columnheaders  # exp_plot: each CSV block starts with a header line
set datafile separator comma
set style fill solid 0.6
set boxwidth 0.6
set ylabel 'bits per pixel'
set yrange [0:*]
set xrange [-0.6:3.6]
set xtics rotate by -15 font ',8'
set rmargin 12
set bmargin 6
set grid ytics
plot 'sizes.csv' using 0:2:xtic(1) with boxes notitle, '' using 0:($2+5):2 with labels notitle
