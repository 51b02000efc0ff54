"""Pictures: feature maps and buffers as images (:mod:`.images`), the mesh coloured by per-vertex
values from standard views (:mod:`.render`, :mod:`.surface_plot`: ``uvfeat.plot``), principal
directions drawn as a line field (:mod:`.line_field`), and the interactive viewer
(:mod:`.viewer`, :mod:`.viewer_panel`: ``uvfeat.view``)."""
