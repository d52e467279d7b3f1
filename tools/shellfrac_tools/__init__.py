"""shellfrac's Python tools, as one package: what the command-line scripts in tools/ and the tests share.

Modules:
  cli            fail(): the one way a script stops on bad input (its name, the message, exit 1)
  tables         history, crack and fragment CSV tables read by column name (a partial last line left out)
  results_files  the files of an Exodus result: one file or a complete per-rank set, names taken literally
  exodus         one reader of shellfrac's Exodus results files (netCDF4): coordinates, blocks, variables
  decks          deck text: parameter lines, checked substitutions
  launch         running shellfrac (or any program) serially or under mpiexec, with the environment MPI needs

The scripts in tools/ import it from their own directory; tests put tools/ on sys.path (or PYTHONPATH).
Needs numpy; `exodus` needs netCDF4 (Debian: python3-numpy, python3-netcdf4; /usr/bin/python3 has both).
"""
