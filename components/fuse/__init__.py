"""The support fuse: a load-reduction device between a supported point and the structure, which breaks at a load."""
