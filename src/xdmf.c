#include <config.h>

#include "xdmf.h"

#include <errno.h>
#include <string.h>
#include <unistd.h>

void mimas_xdmf_path(const char *h5path, const char *suffix, char *out, size_t len)
{
    size_t n = strlen(h5path);
    if (n > 3 && !strcmp(h5path + n - 3, ".h5"))
        n -= 3;
    snprintf(out, len, "%.*s%s.xdmf", (int)n, h5path, suffix ? suffix : "");
}

/* Text as an XML attribute value or element content. */
static void xml_text(FILE *fp, const char *s)
{
    for (; *s; s++) {
        switch (*s) {
        case '&': fputs("&amp;", fp); break;
        case '<': fputs("&lt;", fp); break;
        case '>': fputs("&gt;", fp); break;
        case '"': fputs("&quot;", fp); break;
        default: fputc(*s, fp);
        }
    }
}

int xdmf_begin(xdmf_writer *x, const char *path, const char *h5path, mimas_error *err)
{
    memset(x, 0, sizeof *x);
    snprintf(x->path, sizeof x->path, "%s", path);
    snprintf(x->tmp, sizeof x->tmp, "%s.tmp%ld", path, (long)getpid());
    /* the sidecar sits beside the HDF5 file and names it without a folder */
    const char *base = strrchr(h5path, '/');
    snprintf(x->h5name, sizeof x->h5name, "%s", base ? base + 1 : h5path);
    x->fp = fopen(x->tmp, "w");
    if (!x->fp)
        return mimas_error_set(err, MIMAS_EIO, "%s: cannot write: %s", path, strerror(errno));
    fputs("<?xml version=\"1.0\" ?>\n<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n"
          "<Xdmf xmlns:xi=\"http://www.w3.org/2001/XInclude\" Version=\"2.0\">\n <Domain>\n",
          x->fp);
    return MIMAS_OK;
}

int xdmf_end(xdmf_writer *x, int ok, mimas_error *err)
{
    if (!x->fp)
        return MIMAS_OK;
    if (ok)
        fputs(" </Domain>\n</Xdmf>\n", x->fp);
    int bad = ferror(x->fp) != 0;
    bad |= fclose(x->fp) != 0;
    x->fp = NULL;
    if (ok && !bad && rename(x->tmp, x->path) == 0)
        return MIMAS_OK;
    remove(x->tmp);
    return ok ? mimas_error_set(err, MIMAS_EIO, "%s: cannot write the XDMF file", x->path)
              : MIMAS_OK;
}

void xdmf_item_whole(xdmf_item *it, const char *dataset, int is_float, int precision, int rank,
                     const unsigned long long *dims)
{
    memset(it, 0, sizeof *it);
    it->dataset = dataset;
    it->is_float = is_float;
    it->precision = precision;
    it->rank = rank;
    it->out_rank = rank;
    for (int d = 0; d < rank; d++)
        it->dims[d] = it->out[d] = it->count[d] = dims[d];
}

void xdmf_item_frame(xdmf_item *it, unsigned long long k, unsigned long long n1)
{
    it->slab = 1;
    it->start[0] = k;
    it->count[0] = 1;
    if (n1 && it->rank > 1)
        it->count[1] = n1;
    it->out_rank = it->rank - 1;
    for (int d = 1; d < it->rank; d++)
        it->out[d - 1] = it->count[d];
}

static void indent_to(FILE *fp, int indent)
{
    fprintf(fp, "%*s", indent, "");
}

static void dims_text(FILE *fp, int rank, const unsigned long long *dims)
{
    for (int d = 0; d < rank; d++)
        fprintf(fp, "%s%llu", d ? " " : "", dims[d]);
}

/* The dataset, read as rank x dims values (a whole dataset may be read in
 * another shape of the same size). */
static void write_source(xdmf_writer *x, int indent, const xdmf_item *it, int rank,
                         const unsigned long long *dims)
{
    indent_to(x->fp, indent);
    fputs("<DataItem Dimensions=\"", x->fp);
    dims_text(x->fp, rank, dims);
    fprintf(x->fp, "\" NumberType=\"%s\" Precision=\"%d\" Format=\"HDF\">",
            it->is_float ? "Float" : "Int", it->precision);
    xml_text(x->fp, x->h5name);
    fputc(':', x->fp);
    xml_text(x->fp, it->dataset);
    fputs("</DataItem>\n", x->fp);
}

void xdmf_write_item(xdmf_writer *x, int indent, const xdmf_item *it)
{
    if (!it->slab) {
        write_source(x, indent, it, it->out_rank, it->out);
        return;
    }
    FILE *fp = x->fp;
    indent_to(fp, indent);
    fputs("<DataItem ItemType=\"HyperSlab\" Dimensions=\"", fp);
    dims_text(fp, it->out_rank, it->out);
    fputs("\">\n", fp);
    /* start, stride and count, one row each */
    indent_to(fp, indent + 1);
    fprintf(fp, "<DataItem Dimensions=\"3 %d\" Format=\"XML\">", it->rank);
    for (int d = 0; d < it->rank; d++)
        fprintf(fp, " %llu", it->start[d]);
    for (int d = 0; d < it->rank; d++)
        fputs(" 1", fp);
    for (int d = 0; d < it->rank; d++)
        fprintf(fp, " %llu", it->count[d]);
    fputs(" </DataItem>\n", fp);
    write_source(x, indent + 1, it, it->rank, it->dims);
    indent_to(fp, indent);
    fputs("</DataItem>\n", fp);
}

void xdmf_item_shape(xdmf_item *it, int rank, const unsigned long long *out)
{
    it->out_rank = rank;
    for (int d = 0; d < rank; d++)
        it->out[d] = out[d];
}

static void attribute_open(xdmf_writer *x, int indent, const char *name, const char *type,
                           const char *center)
{
    indent_to(x->fp, indent);
    fputs("<Attribute Name=\"", x->fp);
    xml_text(x->fp, name);
    fprintf(x->fp, "\" AttributeType=\"%s\" Center=\"%s\">\n", type, center);
}

static void attribute_close(xdmf_writer *x, int indent)
{
    indent_to(x->fp, indent);
    fputs("</Attribute>\n", x->fp);
}

void xdmf_write_attribute(xdmf_writer *x, int indent, const char *name, const char *type,
                          const char *center, const xdmf_item *it)
{
    attribute_open(x, indent, name, type, center);
    xdmf_write_item(x, indent + 1, it);
    attribute_close(x, indent);
}

void xdmf_write_joined(xdmf_writer *x, int indent, const char *name, const char *type,
                       const char *center, const xdmf_item *items, int n)
{
    FILE *fp = x->fp;
    attribute_open(x, indent, name, type, center);
    indent_to(fp, indent + 1);
    fputs("<DataItem ItemType=\"Function\" Function=\"JOIN(", fp);
    for (int k = 0; k < n; k++)
        fprintf(fp, "%s$%d", k ? ", " : "", k);
    fputs(")\" Dimensions=\"", fp);
    dims_text(fp, items[0].out_rank, items[0].out);
    fprintf(fp, " %d\">\n", n);
    for (int k = 0; k < n; k++)
        xdmf_write_item(x, indent + 2, &items[k]);
    indent_to(fp, indent + 1);
    fputs("</DataItem>\n", fp);
    attribute_close(x, indent);
}
