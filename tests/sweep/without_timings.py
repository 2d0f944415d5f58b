"""Prints a sweep's results.csv without its timing columns (seconds, wall_seconds): what two
engines that ran the same jobs must agree on. Usage: without_timings.py results.csv"""
import csv
import sys

rows = list(csv.reader(open(sys.argv[1], newline="")))
keep = [i for i, name in enumerate(rows[0]) if name not in ("seconds", "wall_seconds")]
for row in rows:
    print(",".join(row[i] for i in keep))
