"""
description: robot descriptions in and out, one reader and one writer per format, one model for
all: files to the frozen model with source locations, and text edits back on the original bytes.
Nothing above this layer imports a format's folder (an import-linter contract): the layers
above reach the formats through the format-neutral modules.

- format-neutral: ``loader`` (``load(path)``: a file to its format's reader, by content; what
  the include graph, ``-o`` and stdin need), ``model`` (the frozen dataclasses: Robot, Link,
  Joint, Inertial, ... each with its ``Source``), ``writing`` (how values are written, in
  each format's words), ``placement`` (a link's new values to its format's writer's edits),
  ``editing`` (the texts a fix may touch), ``edits`` (text edits on the original bytes, and
  atomic writes, through symbolic links; stale temporary files of killed writes removed; our
  writers one at a time), ``reads`` (what a load read, so that an edit is written only on the
  text it was computed on), ``overlay`` (the texts ``--fix``'s passes read), ``xmlparse``,
  ``safexml``, ``xmlspan``, ``lines`` (XML read as the parsers do, within bounds; where an
  element stands in the text; lines as XML counts them), ``output_paths`` (a named output file
  never through a symbolic link), ``xacro_limits`` (the bounds of a macro expansion),
  ``package_files`` (bounded file checks), ``redaction`` (what the environment gave an
  expansion, kept out of what is printed: ``--redact-env``).
- ``urdf/``: URDF and xacro (the reader, the real xacro in a bounded sandbox, ``$(find)`` and
  ``package://`` without ROS, the ``<inertial>`` block, and ``placement/``: values written as a
  xacro author would).
- ``mjcf/``: MJCF, as MuJoCo's compiler reads it, and its ``<inertial>`` writer.
"""
