"""The elastic-plastic contact laws (Yigit–Christoforou, Stronge, the FE-calibrated epp) and the first yield they share."""
