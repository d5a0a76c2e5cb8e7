"""The inspector: canonical traces read back (``trace``) and the one offline page that replays
them against the supervisors (``page``)."""
