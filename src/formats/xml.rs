//! A tiny element tree rendered through quick-xml, shared by the XML writers (SDFormat, MJCF,
//! package.xml). Text and attribute values are escaped by quick-xml.

use quick_xml::Writer;
use quick_xml::events::{BytesDecl, BytesText, Event};

/// An XML element with attributes, text and children.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct El {
    name: String,
    attrs: Vec<(String, String)>,
    text: Option<String>,
    children: Vec<El>,
}

impl El {
    /// An element called `name`.
    pub fn new(name: &str) -> El {
        El {
            name: name.to_string(),
            ..El::default()
        }
    }

    /// Adds an attribute.
    pub fn attr(mut self, key: &str, value: impl ToString) -> El {
        self.attrs.push((key.to_string(), value.to_string()));
        self
    }

    /// Sets the text content.
    pub fn text(mut self, text: impl ToString) -> El {
        self.text = Some(text.to_string());
        self
    }

    /// Adds a child.
    pub fn child(mut self, child: El) -> El {
        self.children.push(child);
        self
    }

    /// Adds a child in place.
    pub fn push(&mut self, child: El) {
        self.children.push(child);
    }

    /// Adds children.
    pub fn children(mut self, children: impl IntoIterator<Item = El>) -> El {
        self.children.extend(children);
        self
    }

    /// Shorthand for `<name>text</name>`.
    pub fn leaf(name: &str, text: impl ToString) -> El {
        El::new(name).text(text)
    }

    fn write(&self, w: &mut Writer<Vec<u8>>) -> std::io::Result<()> {
        let mut el = w.create_element(self.name.as_str());
        for (k, v) in &self.attrs {
            el = el.with_attribute((k.as_str(), v.as_str()));
        }
        match (&self.text, self.children.is_empty()) {
            (None, true) => {
                el.write_empty()?;
            }
            (Some(t), true) => {
                el.write_text_content(BytesText::new(t))?;
            }
            (text, false) => {
                el.write_inner_content(|w| {
                    if let Some(t) = text {
                        w.write_event(Event::Text(BytesText::new(t)))?;
                    }
                    for c in &self.children {
                        c.write(w)?;
                    }
                    Ok(())
                })?;
            }
        }
        Ok(())
    }

    /// The document text with an XML declaration, two-space indentation and a final newline.
    pub fn to_document(&self) -> String {
        let mut w = Writer::new_with_indent(Vec::new(), b' ', 2);
        // Writing into a Vec cannot fail.
        let _ = w.write_event(Event::Decl(BytesDecl::new("1.0", Some("utf-8"), None)));
        let _ = self.write(&mut w);
        let mut s = String::from_utf8(w.into_inner()).unwrap_or_default();
        s.push('\n');
        s
    }
}

/// Space-separated numbers, shortest round-trip form.
pub fn nums(values: &[f64]) -> String {
    values
        .iter()
        .map(|v| fmt_num(*v))
        .collect::<Vec<_>>()
        .join(" ")
}

/// A number in its shortest round-trip form, with `-0` written as `0`.
pub fn fmt_num(v: f64) -> String {
    if v == 0.0 {
        "0".to_string()
    } else {
        format!("{v}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn escapes_text_and_attributes() {
        let doc = El::new("a")
            .attr("name", "x\"<y>")
            .child(El::leaf("b", "1 < 2 & 3"))
            .to_document();
        assert!(doc.contains("&lt;"));
        assert!(doc.contains("&amp;"));
        assert!(doc.contains("name=\"x&quot;&lt;y&gt;\""));
    }
}
