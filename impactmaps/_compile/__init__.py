"""numba's compile and cache plumbing, beneath every layer: kernels compiled on first use, a helper process compiling beside the first run, the background warm-up."""
