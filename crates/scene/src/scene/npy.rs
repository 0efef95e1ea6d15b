//! The header of a `.npy` file, read as numpy reads it: a Python dict
//! literal with the keys `descr`, `fortran_order` and `shape`, in any
//! order, with any spacing, either quote style and trailing commas
//! (`{'descr': '<f8', 'fortran_order': False, 'shape': (3, 4), }` and
//! `{"shape":(3,4),"fortran_order":True,"descr":"<f4"}` alike).

/// What a `.npy` header says about the array after it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(super) struct NpyHeader {
    /// The values' type as numpy writes it (`<f8`, `>f4`, ...).
    pub descr: String,
    /// Whether the values are stored column by column (Fortran order).
    pub fortran_order: bool,
    /// The array's extent along each axis.
    pub shape: Vec<usize>,
}

/// A value of the header's dict.
enum Value {
    Str(String),
    Bool(bool),
    Tuple(Vec<usize>),
}

/// A cursor over the header's text.
struct Cursor<'a> {
    text: &'a str,
    at: usize,
}

impl Cursor<'_> {
    /// The next character after blanks, not taken.
    fn peek(&mut self) -> Option<char> {
        let rest = &self.text[self.at..];
        self.at += rest.len() - rest.trim_start().len();
        self.text[self.at..].chars().next()
    }

    /// Takes `c` (after blanks), or says what stands in its place.
    fn expect(&mut self, c: char) -> Result<(), String> {
        match self.peek() {
            Some(found) if found == c => {
                self.at += c.len_utf8();
                Ok(())
            }
            found => Err(format!("expected '{c}' at {}", self.found(found))),
        }
    }

    /// Takes `c` (after blanks) if it is next.
    fn take(&mut self, c: char) -> bool {
        let next = self.peek() == Some(c);
        if next {
            self.at += c.len_utf8();
        }
        next
    }

    /// Where the cursor stands, as a message names it.
    fn found(&self, c: Option<char>) -> String {
        match c {
            Some(c) => format!("character {} ('{}')", self.at, c.escape_default()),
            None => "the header's end".to_string(),
        }
    }

    /// A quoted string, either quote style, without escapes.
    fn string(&mut self) -> Result<String, String> {
        let quote = match self.peek() {
            Some(q @ ('\'' | '"')) => q,
            c => return Err(format!("expected a quoted string at {}", self.found(c))),
        };
        let start = self.at + 1;
        let len = self.text[start..]
            .find(quote)
            .ok_or("a string is not closed")?;
        self.at = start + len + 1;
        Ok(self.text[start..start + len].to_string())
    }

    /// A word of letters and digits (`True`, `False`, `3`, `3L`).
    fn word(&mut self) -> &str {
        self.peek();
        let rest = &self.text[self.at..];
        let len = rest
            .find(|c: char| !c.is_ascii_alphanumeric() && c != '_')
            .unwrap_or(rest.len());
        self.at += len;
        &rest[..len]
    }

    /// A tuple of counts: `()`, `(3,)`, `(3, 4)`, `(3, 4,)`.
    fn tuple(&mut self) -> Result<Vec<usize>, String> {
        self.expect('(')?;
        let mut dims = Vec::new();
        while !self.take(')') {
            let word = self.word();
            // Python 2's numpy wrote long integers as `3L`.
            let digits = word.strip_suffix('L').unwrap_or(word);
            let dim = digits
                .parse::<usize>()
                .map_err(|_| format!("the shape holds {word:?}, not a count"))?;
            dims.push(dim);
            if !self.take(',') {
                self.expect(')')?;
                break;
            }
        }
        Ok(dims)
    }

    /// A value: a string, `True`/`False` or a tuple.
    fn value(&mut self) -> Result<Value, String> {
        match self.peek() {
            Some('\'' | '"') => self.string().map(Value::Str),
            Some('(') => self.tuple().map(Value::Tuple),
            c => match self.word() {
                "True" => Ok(Value::Bool(true)),
                "False" => Ok(Value::Bool(false)),
                _ => Err(format!(
                    "expected a string, True, False or a tuple at {}",
                    self.found(c)
                )),
            },
        }
    }
}

/// The header `text` read, or what is wrong with it, in numpy's terms.
pub(super) fn parse_header(text: &str) -> Result<NpyHeader, String> {
    let mut c = Cursor { text, at: 0 };
    c.expect('{')?;
    let (mut descr, mut fortran_order, mut shape) = (None, None, None);
    while !c.take('}') {
        let key = c.string()?;
        if !matches!(key.as_str(), "descr" | "fortran_order" | "shape") {
            let shown: String = key.chars().take(20).collect();
            return Err(format!(
                "the header has a key {shown:?} numpy does not write"
            ));
        }
        c.expect(':')?;
        let value = c.value()?;
        let slot_taken = match (key.as_str(), value) {
            ("descr", Value::Str(s)) => descr.replace(s).is_some(),
            ("fortran_order", Value::Bool(b)) => fortran_order.replace(b).is_some(),
            ("shape", Value::Tuple(t)) => shape.replace(t).is_some(),
            _ => return Err(format!("the header's '{key}' has the wrong type")),
        };
        if slot_taken {
            return Err(format!("the header gives '{key}' twice"));
        }
        if !c.take(',') {
            c.expect('}')?;
            break;
        }
    }
    if let Some(rest) = Some(c.text[c.at..].trim()).filter(|r| !r.is_empty()) {
        let shown: String = rest.chars().take(20).collect();
        return Err(format!("the header goes on after its dict ({shown:?})"));
    }
    let missing = |k: &str| format!("the header has no '{k}'");
    Ok(NpyHeader {
        descr: descr.ok_or_else(|| missing("descr"))?,
        fortran_order: fortran_order.ok_or_else(|| missing("fortran_order"))?,
        shape: shape.ok_or_else(|| missing("shape"))?,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn header(descr: &str, fortran_order: bool, shape: &[usize]) -> NpyHeader {
        NpyHeader {
            descr: descr.to_string(),
            fortran_order,
            shape: shape.to_vec(),
        }
    }

    #[test]
    fn numpy_s_own_header_is_read() {
        let h = "{'descr': '<f8', 'fortran_order': False, 'shape': (3, 4), }          \n";
        assert_eq!(parse_header(h), Ok(header("<f8", false, &[3, 4])));
    }

    #[test]
    fn any_spacing_quotes_order_and_trailing_commas_are_read() {
        for (h, want) in [
            (
                "{'descr':'<f8','fortran_order':True,'shape':(3,4)}",
                header("<f8", true, &[3, 4]),
            ),
            (
                "{\"shape\" : ( 3 , 4 , ) , \"fortran_order\" :True, \"descr\":\"<f4\",}",
                header("<f4", true, &[3, 4]),
            ),
            (
                "{ 'fortran_order' : False ,\n 'descr' : '>f8' , 'shape' : (5,) }\n",
                header(">f8", false, &[5]),
            ),
            (
                "{'descr': '<f8', 'fortran_order': False, 'shape': (2L, 3L), }",
                header("<f8", false, &[2, 3]),
            ),
            (
                "{'descr': '<f8', 'fortran_order': False, 'shape': (), }",
                header("<f8", false, &[]),
            ),
        ] {
            assert_eq!(parse_header(h), Ok(want), "{h}");
        }
    }

    #[test]
    fn a_bad_header_is_refused_saying_why() {
        for (h, why) in [
            ("{'descr': '<f8', 'shape': (3, 4)}", "no 'fortran_order'"),
            (
                "{'descr': '<f8', 'fortran_order': 1, 'shape': (3, 4)}",
                "expected a string, True, False",
            ),
            (
                "{'descr': '<f8', 'fortran_order': False, 'shape': (3, -4)}",
                "not a count",
            ),
            (
                "{'descr': '<f8', 'fortran_order': False, 'shape': (3, 4), 'x': 1}",
                "numpy does not write",
            ),
            (
                "{'descr': '<f8', 'descr': '<f4', 'fortran_order': False, 'shape': (3,)}",
                "twice",
            ),
            (
                "{'descr': '<f8', 'fortran_order': False, 'shape': (3, 4)",
                "end",
            ),
            ("{'descr': '<f8, 'fortran_order': False}", "expected '}'"),
            (
                "{'descr': '<f8', 'fortran_order': 'no', 'shape': (3,)}",
                "wrong type",
            ),
            (
                "{'descr': '<f8', 'fortran_order': False, 'shape': (3,)} x",
                "goes on",
            ),
        ] {
            let e = parse_header(h).unwrap_err();
            assert!(e.contains(why), "{h}: {e}");
        }
    }
}
