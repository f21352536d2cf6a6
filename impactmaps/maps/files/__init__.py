"""Map files: packed arrays, the resumable store and its lock, shipped results."""
