"""The compiler pipeline in one call: load -> validate -> canonicalise -> tables -> image."""

import os
from dataclasses import dataclass

from .canonical import canonicalise
from .errors import InputError
from .image import pack
from .load_automata import load_automata
from .load_supervisor import load_supervisor
from .model import Model
from .naming import model_identifier
from .tables import Tables, build_tables


@dataclass(frozen=True)
class Compiled:
    name: str          # identifier-safe model name, used for generated file names
    model: Model
    tables: Tables
    image: bytes


def load(paths):
    """One supervisor.yaml, or one or more Nadzoru 2 XML automata (one local supervisor each)."""
    paths = list(paths)
    xml = [p for p in paths if p.lower().endswith(".xml")]
    if xml and len(xml) != len(paths):
        raise InputError(paths[0], "", "give either one supervisor.yaml or XML automata, not both")
    if not xml and len(paths) != 1:
        raise InputError(paths[1], "", "a compiled supervisor is one file; give one .yaml at a time")
    return load_automata(paths) if xml else load_supervisor(paths[0])


def model_name(paths, name=None):
    """The model's name: ``name`` if given, else the first input's file stem, as an identifier
    (naming.model_identifier)."""
    return model_identifier(name or os.path.splitext(os.path.basename(paths[0]))[0], paths[0])


def compile_inputs(paths, name=None, names=True):
    """Run the whole pipeline; raises InputError on bad input."""
    return compile_spec(load(paths), paths, name, names)


def compile_spec(spec, paths, name=None, names=True):
    """The pipeline after loading: canonicalise, build tables, pack the image."""
    model = canonicalise(spec)
    tables = build_tables(model)
    return Compiled(model_name(paths, name), model, tables, pack(tables, spec.source, names=names))
