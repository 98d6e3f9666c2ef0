"""KanjiVG characters, demonstrations and training batches."""
