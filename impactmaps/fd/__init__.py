"""Finite-difference Rayleigh beam with a layered elastic-plastic cross-section."""
