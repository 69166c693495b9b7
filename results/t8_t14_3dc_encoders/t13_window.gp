set key noenhanced  # exp_plot: titles are plain names
set xlabel 'window half-width (codes)'
set ylabel 'blocks at the exact optimum (%)'
set y2label 'error left vs optimum (% of sum dN^2)'
set ytics nomirror
set y2tics
set grid
set key center right
plot 't13_window.dat' using 1:2 with linespoints lw 2 title 'at optimum (common base)', '' using 1:3 axes x1y2 with linespoints lw 2 title 'error left (common base)', '' using 1:5 with linespoints lw 2 dt 2 title 'at optimum (fast base)', '' using 1:6 axes x1y2 with linespoints lw 2 dt 2 title 'error left (fast base)'

