// placeholder: report.html is being written
