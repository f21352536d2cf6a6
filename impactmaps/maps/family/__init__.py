"""What a map is: the families, their layouts and registry, statuses, regimes, structures and the refinement tree."""
