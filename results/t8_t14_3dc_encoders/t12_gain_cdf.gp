set key noenhanced  # exp_plot: titles are plain names
set xlabel 'per-block error reduction of the optimal encoder over common (% of sum dN^2)'
set ylabel 'fraction of blocks'
set grid
set key bottom right
set logscale x
set xrange [0.01:100]
plot for [i=0:3] 't12_gain_cdf.dat' index i using ($1>0.01?$1:0.01):2 with steps lw 2 title word('bumps ridges noise hood', i+1)

