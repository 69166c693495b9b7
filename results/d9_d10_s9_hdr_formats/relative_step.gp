set datafile separator comma
set logscale xy
set grid
set format x '10^{%L}'
set format y '10^{%L}'
set xlabel 'stored value'
set ylabel 'quantisation step / value'
set yrange [1e-4:10]
set key bottom left
plot for [i=2:6] 'relative_step.csv' using 1:i with lines lw 2 title columnheader(i)
