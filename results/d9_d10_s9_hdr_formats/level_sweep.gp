set key noenhanced  # exp_plot: titles are plain names
set datafile columnheaders  # exp_plot: each CSV block starts with a header line
set datafile separator comma
set logscale x
set grid
set format x '10^{%L}'
set xlabel 'absolute level of the interior scene (x 1)'
set ylabel 'mean display-code error'
set key outside right
set logscale y
set yrange [1e-3:200]
plot 'level_sweep.csv' using 1:($5+1e-3) with lines lw 2 title 'R11G11B10F, no scaling', '' using 1:($6+1e-3) with lines lw 2 title 'R11G11B10F, c/l', '' using 1:($8+1e-3) with lines lw 2 title 'RGBM, no scaling', '' using 1:($10+1e-3) with lines lw 2 title 'RGBM, window', '' using 1:($3+1e-3) with lines dt 2 title 'RGBA16F, c/l', '' using 1:($13+1e-3) with lines dt 3 title 'RGB10 0..2, window'
