"""Moving users' existing projects onto swarmvm: edits of their own files, as the docs describe
(``switch``: an OpenSwarm ARGoS project's build files and includes onto the C++ drop-in)."""
