"""The Python runtime: standalone, standard-library-only modules that generated Python and
Pi-puck targets receive as copies, and that the compiler imports as swarmvm.runtime_py.*."""
