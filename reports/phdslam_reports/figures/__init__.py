"""One module per figure family; each returns a matplotlib Figure or None when data are missing."""
