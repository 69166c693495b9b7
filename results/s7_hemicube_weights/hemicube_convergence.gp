set key noenhanced  # exp_plot: titles are plain names
set datafile separator comma
set logscale xy
set grid
set xlabel 'texels per hemicube face side'
set ylabel '|sum of centre-cosine weights / pi - 1|'
plot 'hemicube_convergence.csv' every ::1 using 1:2 with linespoints pt 7 title 'centre-cosine weights'

