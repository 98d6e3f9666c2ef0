"""Planning: the policy loop, the slot batcher, stroke ordering and ``plan``."""
