"""Package data: the Jinja templates of every target, one folder per target (read through
importlib.resources by swarmvm.compiler.render; nothing here is imported as code)."""
