"""
lint: rules over the analysed robot, and findings out.

``runner`` loads each file, analyses it once and runs every enabled rule of the ``catalog``
(the one registry of ``rules/``, one module per rule; the contract is in
:mod:`inertia_kit.lint.rules`), with their typed ``options``, the ``config`` (and
``config_files``) and the ``suppress`` comments, whose use ``unused`` judges (IN090);
``add_noqa`` writes a comment for every finding (placed by ``markup``); ``repository_links``
refuses to write a robot file that links out of its repository; ``merge`` joins the results of
several files; ``scan`` (``scan_pool``, ``scan_record``, ``scan_summary``) lints an asset
library one asset at a time under limits, into a resumable JSON Lines record (``inertia-kit
scan``), ``scan_dask`` on a Dask cluster (``--dask``);
``output/`` prints them, one module per format; ``documents`` finds each rule's document.
"""
