set key noenhanced  # exp_plot: titles are plain names
set datafile separator comma
set xlabel 'distance of the light to the wall (m), radius 5 m'
set ylabel 'light in the next room / light in its own room'
set y2label 'light-volume pixels rejected by the clip volume'
set y2tics
set ytics nomirror
set key top right
set grid
plot 'leak_vs_distance.csv' every ::1 using 1:2 with linespoints pt 7 title 'leak, unshadowed', '' every ::1 using 1:3 with linespoints pt 6 title 'leak, with clip volume', '' every ::1 using 1:4 axes x1y2 with lines dt 2 title 'pixels rejected (right axis)'

