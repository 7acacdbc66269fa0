"""Study drivers: which runs a document needs, in which batches, and how they combine."""
