"""A node that never starts: it fails as it is imported."""

raise RuntimeError("this student's node is broken")
