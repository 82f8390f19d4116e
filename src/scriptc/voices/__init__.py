"""Voice backends: synthesise lines into clips with word timings."""
