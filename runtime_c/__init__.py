"""Package data: the C runtime (C99), copied into generated C, Kilobot and CapBot targets."""
