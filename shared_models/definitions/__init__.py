"""Interface definition files (``.msg``, ``.srv``, ``.action``) as Skydeck types.

    parser.py    the files' text -> plain data (ROS 1's syntax and ROS 2's)
    builder.py   plain data -> message and service classes, the same kind as shared_models' own
    actions.py   an action's classes, and the ones ROS 2 and ROS 1's actionlib derive from it
    index.py     where packages are on disk: shipped (shared_models/packages/) and workspaces
    loader.py    a package's files loaded in dependency order; definitions sent to, and learned
                 from, another process (how the core learns a node's types)
    errors.py    DefinitionError (file and line), DefinitionConflict

See docs/ros.md, "Custom interfaces".
"""
