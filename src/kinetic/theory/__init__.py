"""Theory curves: one module per document (``visco2008``, ``montanero2007``, ...)."""
