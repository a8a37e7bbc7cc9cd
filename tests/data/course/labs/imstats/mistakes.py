"""Lab 13's mistakes table: each case is the reference with one function redefined, the
exercise it must lose points in, and the words its diagnosis must contain."""

MISTAKES = {
    "normalised histogram": ("lab13.ex1", """
        def histogram(image, bins=256):
            counts = np.bincount(np.asarray(image).astype(np.int64).ravel() * bins // 256, minlength=bins)
            return counts / counts.sum()
        """, ["normalised"]),
    "np.histogram over the image's own range": ("lab13.ex1", """
        def histogram(image, bins=256):
            return np.histogram(image, bins)[0]
        """, ["own darkest and brightest"]),
    "cumulative histogram": ("lab13.ex1", """
        def histogram(image, bins=256):
            return np.cumsum(np.bincount(np.asarray(image).astype(np.int64).ravel() * bins // 256,
                                         minlength=bins))
        """, ["cumulative"]),
    "bins ignored": ("lab13.ex1", """
        def histogram(image, bins=256):
            return np.bincount(np.asarray(image).ravel(), minlength=256)
        """, ["histogram(image, bins=16)"]),
    "counts in a float array": ("lab13.ex1", """
        def histogram(image, bins=256):
            counts = np.zeros(bins)
            np.add.at(counts, np.asarray(image).astype(np.int64).ravel() * bins // 256, 1)
            return counts
        """, ["has dtype float64", "must be integer"]),
    "stretch in uint8": ("lab13.ex2", """
        def stretch(image):
            low, high = image.min(), image.max()
            if high == low:
                return np.zeros_like(image)
            return (image - low) * np.uint8(255) // (high - low)
        """, ["uint8", "wraps around"]),
    "stretch truncated": ("lab13.ex2", """
        def stretch(image):
            image = np.asarray(image, float)
            low, high = image.min(), image.max()
            if high == low:
                return np.zeros(image.shape, np.uint8)
            return ((image - low) * 255.0 / (high - low)).astype(np.uint8)
        """, ["truncated"]),
    "stretch without subtracting the minimum": ("lab13.ex2", """
        def stretch(image):
            image = np.asarray(image, float)
            return np.round(image * 255.0 / image.max()).astype(np.uint8)
        """, ["minimum is not subtracted"]),
    "stretch to 0..1": ("lab13.ex2", """
        def stretch(image):
            image = np.asarray(image, float)
            low, high = image.min(), image.max()
            return (image - low) / (high - low) if high > low else np.zeros(image.shape)
        """, ["0..1"]),
    "stretch of a constant image divides by zero": ("lab13.ex2", """
        def stretch(image):
            image = np.asarray(image, float)
            low, high = image.min(), image.max()
            return np.round(np.nan_to_num((image - low) * 255.0 / (high - low))).astype(np.uint8) \\
                if high > low else np.full(image.shape, 255, np.uint8)
        """, ["stretch(constant image) differs"]),
    "stretch returns float64": ("lab13.ex2", """
        def stretch(image):
            image = np.asarray(image, float)
            low, high = image.min(), image.max()
            if high == low:
                return np.zeros(image.shape)
            return np.round((image - low) * 255.0 / (high - low))
        """, ["dtype float64"]),
}
