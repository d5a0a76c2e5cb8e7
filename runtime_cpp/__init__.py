"""Package data: the header-only C++17 runtime, copied into generated ARGoS targets."""
