"""Course content: locating a course, loading chapters and exercises, drawing variants."""
