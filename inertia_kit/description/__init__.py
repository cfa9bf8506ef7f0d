"""
description: robot descriptions in and out: files to the frozen model with source locations,
and text edits back on the original bytes.

- ``loader``: ``load(path)`` (``xmlparse`` reads the bytes as the URDF parsers do, ``safexml``
  bounds and secures the parse, ``builder`` makes the model); ``xacro_expand`` (with
  ``xacro_session``, the hooks in xacro, ``xacro_source_map`` and ``xacro_errors``): xacro
  through the real package, with a source map, within the time, memory and element limits of
  ``xacro_limits`` (in a forked child process: ``xacro_sandbox``; YAML through
  ``xacro.load_yaml`` bounded by ``xacro_yaml``); ``xacro_detect``: whether
  a file is xacro, without importing any of that;
  ``packages``: ``$(find)`` and ``package://`` without ROS (finding packages:
  ``package_lookup``; file checks, ``package.xml`` names and bounded walks: ``package_files``).
- ``model``: the frozen dataclasses (Robot, Link, Joint, Inertial, ... each with its ``Source``).
- ``inertial_xml``: an ``<inertial>`` block as text; ``xmlspan``: where an element stands in the
  original text; ``lines``: lines as XML counts them (a lone CR ends one), in one place;
  ``edits``: text edits on the original bytes, and atomic writes (through
  symbolic links; stale temporary files of killed writes removed; our writers one at a time);
  ``reads``: what a load read (a digest of each file), so that an edit is written only on the
  text it was computed on; ``output_paths``: a named output file never through a symbolic link.
- ``redaction``: what the environment gave a xacro expansion, kept out of what is printed
  (``--redact-env``).
"""
