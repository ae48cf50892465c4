"""Figures, tables and an HTML report built from phdslam results folders.

The package reads only the files a ``phdslam run --out DIR`` invocation writes (see
``validation/README.md``); it never runs an estimator.
"""
