set key noenhanced  # exp_plot: titles are plain names
set datafile columnheaders  # exp_plot: each CSV block starts with a header line
set datafile separator comma
set logscale x
set xlabel 'threshold (deviation of full blur)'
set ylabel 'RMS error'
set grid
set key right center
plot 'threshold_curves.csv' index 0 using 2:4 with linespoints lw 2 title 'pinwheel 4 bilinear', '' index 1 using 2:4 with linespoints title 'diagonal 4 bilinear', '' index 2 using 2:4 with linespoints dt 2 title 'direct 8 point', 0.068633 with lines lc rgb 'black' title 'aliased (no filter)', '' index 0 using 2:3 with linespoints dt 3 title 'pinwheel, all pixels', 0.014171 with lines dt 3 lc rgb 'black' title 'aliased, all pixels'
