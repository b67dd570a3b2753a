/*
 * MpbSpyProbe.java - test_spy.sh's window into a running lcm-spy. lcm-spy
 * instantiates every lcm.spy.SpyPlugin on its class path at start-up; this
 * one, put there with `mpb spy --classpath`, watches lcm-spy's own channel
 * table (what its window shows: channel, type, undecodable count) and the
 * message lcm-spy decoded last on each channel, and prints them:
 *
 *   probe: MPB_STATUS type=daemon_status_t class=mpb.daemon_status_t undecodable=0
 *   probe: MPB_STATUS experiment=spydemo
 *   probe: MPB_STATUS planners[0].name=null
 *
 * each channel's first message (a channel of an unknown type: its type
 * line, class=none), and MPB_STATUS whenever it changes. With
 * MPB_SPY_PROBE_VIEW=CHANNEL it also opens lcm-spy's viewer of that channel
 * (as a double-click would), beside the main window, for the screenshot.
 *
 * lcm-spy adds channels to its map, list and table from its LCM thread, so
 * a snapshot taken meanwhile on the Swing thread can throw (a row the
 * sorter does not know yet). Such a snapshot is taken again 250 ms later
 * ("probe: retry: ..."); "probe: failed: ..." only when 20 in a row fail.
 */
package mpbprobe;

import java.awt.Component;
import java.awt.Container;
import java.awt.Frame;
import java.lang.reflect.Array;
import java.lang.reflect.Field;
import java.lang.reflect.Method;
import java.lang.reflect.Modifier;
import java.util.HashMap;
import java.util.Map;
import javax.swing.Action;
import javax.swing.JDesktopPane;
import javax.swing.JFrame;
import javax.swing.JTable;
import javax.swing.SwingUtilities;

public class MpbSpyProbe implements lcm.spy.SpyPlugin
{
    private final Map<String, String> printed = new HashMap<>();
    private final String view = System.getenv("MPB_SPY_PROBE_VIEW");
    private boolean viewOpen = false;
    private int failedInARow = 0;
    private static final int FAILURES_TOLERATED = 20;

    public MpbSpyProbe()
    {
        Thread t = new Thread(this::watch, "mpb-spy-probe");
        t.setDaemon(true);
        t.start();
    }

    public boolean canHandle(long fingerprint) { return false; }

    public Action getAction(JDesktopPane desktop, lcm.spy.ChannelData cd) { return null; }

    private void watch()
    {
        try {
            JTable table = null;
            while (table == null) {
                Thread.sleep(100);
                table = findTable();
            }
            System.out.println("probe: watching");
            System.out.flush();
            Object spy = spyOf(table);
            final JTable tbl = table;
            while (true) {
                Thread.sleep(250);
                SwingUtilities.invokeAndWait(() -> snapshot(tbl, spy));
            }
        } catch (Exception e) {
            System.out.println("probe: failed: " + e);
            System.out.flush();
        }
    }

    /* The channel table of the frame titled "LCM Spy". */
    private static JTable findTable()
    {
        for (Frame f : Frame.getFrames())
            if ("LCM Spy".equals(f.getTitle())) {
                JTable t = findIn(f);
                if (t != null)
                    return t;
            }
        return null;
    }

    private static JTable findIn(Component c)
    {
        if (c instanceof JTable)
            return (JTable) c;
        if (c instanceof Container)
            for (Component k : ((Container) c).getComponents()) {
                JTable t = findIn(k);
                if (t != null)
                    return t;
            }
        return null;
    }

    private static Object field(Object o, Class<?> cls, String name) throws Exception
    {
        Field f = cls.getDeclaredField(name);
        f.setAccessible(true);
        return f.get(o);
    }

    /* The table's model is a TableSorter over Spy's ChannelTableModel, an
     * inner class whose outer instance is the Spy. */
    private static Object spyOf(JTable table) throws Exception
    {
        Object model = field(table.getModel(), lcm.util.TableSorter.class, "tableModel");
        return field(model, model.getClass(), "this$0");
    }

    private void snapshot(JTable table, Object spy)
    {
        try {
            @SuppressWarnings("unchecked")
            Map<String, lcm.spy.ChannelData> channels =
                (Map<String, lcm.spy.ChannelData>) field(spy, spy.getClass(), "channelMap");
            /* The cells are read from Spy's own model, by the channel's
             * row there: the sorter in front of it re-sorts from the LCM
             * thread, so two cells of one of its rows, read one after the
             * other, may belong to two channels. */
            javax.swing.table.TableModel model = (javax.swing.table.TableModel)
                field(table.getModel(), lcm.util.TableSorter.class, "tableModel");
            for (int row = 0; row < model.getRowCount(); row++) {
                String channel = String.valueOf(model.getValueAt(row, 0));
                lcm.spy.ChannelData cd = channels.get(channel);
                /* A channel of an unknown type has no last message. */
                if (cd == null || (cd.last == null && cd.cls != null))
                    continue;
                if (cd.row != row)
                    throw new IllegalStateException(channel + " at row " + row
                                                    + ", its data says " + cd.row);
                StringBuilder sb = new StringBuilder();
                String p = "probe: " + channel + " ";
                sb.append(p).append("type=").append(model.getValueAt(row, 1))
                  .append(" class=").append(cd.cls == null ? "none" : cd.cls.getName())
                  .append(" undecodable=").append(model.getValueAt(row, 7)).append('\n');
                if (cd.last != null)
                    dump(sb, p, "", cd.last, 0);
                String text = sb.toString();
                String before = printed.get(channel);
                if (before == null || (channel.equals("MPB_STATUS") && !before.equals(text))) {
                    printed.put(channel, text);
                    System.out.print(text);
                    System.out.flush();
                }
                if (channel.equals(view) && !viewOpen)
                    openViewer(spy, cd);
            }
            failedInARow = 0;
        } catch (Exception e) {
            failedInARow++;
            System.out.println((failedInARow < FAILURES_TOLERATED ? "probe: retry: "
                                                                   : "probe: failed: ") + e);
            System.out.flush();
        }
    }

    private void openViewer(Object spy, lcm.spy.ChannelData cd) throws Exception
    {
        Method m = spy.getClass().getDeclaredMethod("createViewer", lcm.spy.ChannelData.class);
        m.setAccessible(true);
        m.invoke(spy, cd);
        JFrame frame = cd.viewerFrame;
        if (frame != null)
            frame.setBounds(800, 0, 650, 600);
        viewOpen = true;
        System.out.println("probe: viewer open " + cd.name);
    }

    /* The public fields of a decoded LCM message, one line each; arrays of
     * messages element by element; long strings cut. */
    private static void dump(StringBuilder sb, String p, String prefix, Object o,
                             int depth) throws Exception
    {
        for (Field f : o.getClass().getFields()) {
            if (Modifier.isStatic(f.getModifiers()))
                continue;
            Object v = f.get(o);
            String name = prefix + f.getName();
            if (v != null && v.getClass().isArray()) {
                int n = Array.getLength(v);
                sb.append(p).append(name).append(".length=").append(n).append('\n');
                for (int i = 0; i < n && i < 8; i++) {
                    Object e = Array.get(v, i);
                    if (e != null && e.getClass().getName().startsWith("mpb.") && depth < 2)
                        dump(sb, p, name + "[" + i + "].", e, depth + 1);
                    else if (e instanceof String)
                        sb.append(p).append(name).append("[").append(i).append("]=")
                          .append(cut((String) e)).append('\n');
                }
            } else if (v != null && v.getClass().getName().startsWith("mpb.") && depth < 2) {
                dump(sb, p, name + ".", v, depth + 1);
            } else {
                sb.append(p).append(name).append('=')
                  .append(v instanceof String ? cut((String) v) : String.valueOf(v))
                  .append('\n');
            }
        }
    }

    private static String cut(String s)
    {
        s = s.replace('\n', ' ');
        return s.length() > 60 ? s.substring(0, 60) + "..." : s;
    }
}
