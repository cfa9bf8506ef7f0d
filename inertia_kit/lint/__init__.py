"""
lint: rules over the analysed robot, and findings out.

``runner`` loads each file, analyses it once and runs every enabled rule of the ``catalog``
(the one registry of ``rules/``, one module per rule; the contract is in
:mod:`inertia_kit.lint.rules`), with their typed ``options``, the ``config`` (and
``config_files``) and the ``suppress`` comments; ``merge`` joins the results of several files;
``output/`` prints them, one module per format; ``documents`` finds each rule's document.
"""
