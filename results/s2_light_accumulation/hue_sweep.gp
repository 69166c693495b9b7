set key noenhanced  # exp_plot: titles are plain names
set datafile separator comma
set xlabel 'hue difference between the two lights (degrees)'
set ylabel 'specular hue error of 4 channels (degrees)'
set key top left
set grid
plot 'hue_sweep.csv' every ::1 using 1:2 with linespoints title 'mean, Phong n=8', '' every ::1 using 1:3 with linespoints title 'max, Phong n=8', '' every ::1 using 1:4 with linespoints title 'mean, Phong n=64', '' every ::1 using 1:5 with linespoints title 'max, Phong n=64'

