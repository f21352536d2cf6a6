"""Plates: the Plate target (Kirchhoff, Mindlin), its Navier, Ritz and static solutions."""
