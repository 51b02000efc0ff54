"""Files uvfeat writes for other tools and for later runs: per-vertex PLY/NPZ and JSON
(:mod:`.writers`), what ``uvfeat compute`` and ``uvfeat batch`` write for one mesh
(:mod:`.feature_files`), textures baked on the mesh's UVs (:mod:`.bake`: ``uvfeat.bake``), and
the warnings of a computation recorded as the notes of their summaries (:mod:`.notes`)."""
