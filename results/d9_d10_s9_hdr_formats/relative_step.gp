set key noenhanced  # exp_plot: titles are plain names
set datafile columnheaders  # exp_plot: each CSV block starts with a header line
set datafile separator comma
set logscale xy
set grid
set format x '10^{%L}'
set format y '10^{%L}'
set xlabel 'stored value'
set ylabel 'quantisation step / value'
set yrange [1e-4:10]
set key bottom left
plot 'relative_step.csv' using 1:2 with lines lw 2 title 'RGBA16F', 'relative_step.csv' using 1:3 with lines lw 2 title 'R11G11B10F', 'relative_step.csv' using 1:4 with lines lw 2 title 'RGBM (RGBA8, range 8)', 'relative_step.csv' using 1:5 with lines lw 2 title 'RGB10 0..2', 'relative_step.csv' using 1:6 with lines lw 2 title 'RGB8 0..1'
