"""Beams: the Beam target and one module per method of its modes and static response."""
